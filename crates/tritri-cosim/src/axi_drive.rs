//! The rust-hdl side of an AXI4 manager port against the Rust memory model
//! ([`tritri_rtl::axi::memory_model`]), for every unit whose port has the
//! `m_axi_` names: the memory's outputs onto the unit's inputs, and the
//! unit's outputs as the memory's [`ManagerSignals`]. Macros, because the
//! units are different types with the same field names.
//!
//! [`ManagerSignals`]: tritri_rtl::axi::memory_model::ManagerSignals

/// Drives `$uut`'s subordinate-side inputs from `$out`
/// (`AxiMemory::outputs()`): OKAY responses, ID 0.
macro_rules! drive_from_memory {
    ($uut:expr, $out:expr, $dw:expr) => {{
        let out = $out;
        $uut.m_axi_arready.next = out.arready;
        $uut.m_axi_rvalid.next = out.rvalid;
        $uut.m_axi_rdata.next = $crate::axi_copy::bits_of::<$dw>(&out.rdata);
        $uut.m_axi_rlast.next = out.rlast;
        $uut.m_axi_rresp.next = 0.into();
        $uut.m_axi_rid.next = false;
        $uut.m_axi_bid.next = false;
        $uut.m_axi_awready.next = out.awready;
        $uut.m_axi_wready.next = out.wready;
        $uut.m_axi_bvalid.next = out.bvalid;
        $uut.m_axi_bresp.next = 0.into();
    }};
}

/// `$uut`'s manager-side outputs, settled, as the memory model reads them.
macro_rules! manager_signals {
    ($uut:expr, $dw:expr) => {
        tritri_rtl::axi::memory_model::ManagerSignals {
            arvalid: $uut.m_axi_arvalid.val(),
            araddr: $uut.m_axi_araddr.val().to_u64(),
            arlen: $uut.m_axi_arlen.val().to_u64(),
            arsize: $uut.m_axi_arsize.val().to_u64(),
            arburst: $uut.m_axi_arburst.val().to_u64(),
            rready: $uut.m_axi_rready.val(),
            awvalid: $uut.m_axi_awvalid.val(),
            awaddr: $uut.m_axi_awaddr.val().to_u64(),
            awlen: $uut.m_axi_awlen.val().to_u64(),
            awsize: $uut.m_axi_awsize.val().to_u64(),
            awburst: $uut.m_axi_awburst.val().to_u64(),
            wvalid: $uut.m_axi_wvalid.val(),
            wdata: $crate::axi_copy::bytes_of::<$dw>($uut.m_axi_wdata.val()),
            wlast: $uut.m_axi_wlast.val(),
            bready: $uut.m_axi_bready.val(),
        }
    };
}

pub(crate) use {drive_from_memory, manager_signals};
